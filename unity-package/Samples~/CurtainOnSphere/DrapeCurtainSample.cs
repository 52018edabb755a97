using UnityEngine;

namespace Drape.Samples.Curtain
{
    /// <summary>Drape sample "Curtain falling on a sphere": add this to an empty GameObject in an empty
    /// scene and press Play. A free 2 m x 2 m cloth falls onto a sphere (Unity SphereCollider,
    /// registered on the cloth) standing on a floor (a plane collider), drapes over it, and falls
    /// asleep once it rests. Every few seconds it is dropped again; the sphere can be moved in the
    /// Scene view while it plays and the cloth reacts (moving a collider wakes it).</summary>
    [AddComponentMenu("Drape/Samples/Curtain On Sphere")]
    public sealed class DrapeCurtainSample : MonoBehaviour
    {
        [Tooltip("Seconds between drops; 0 = drop once.")]
        [Range(0f, 60f)] public float DropEvery = 8f;

        private DrapeCloth _curtain;
        private float _nextDrop;

        private void Start()
        {
            var floor = GameObject.CreatePrimitive(PrimitiveType.Plane);
            floor.name = "Floor";

            var sphere = GameObject.CreatePrimitive(PrimitiveType.Sphere); // radius 0.5 x scale
            sphere.name = "Sphere";
            sphere.transform.position = new Vector3(0f, 0.6f, 0f);
            sphere.transform.localScale = new Vector3(1.2f, 1.2f, 1.2f);

            var curtain = new GameObject("Curtain");
            curtain.SetActive(false);
            // The generated grid lies in local XY hanging down -Y; turned 90 degrees about X it lies
            // flat, 2 m above the floor, centred over the sphere.
            curtain.transform.position = new Vector3(0f, 2f, 1f);
            curtain.transform.rotation = Quaternion.Euler(90f, 0f, 0f);
            curtain.AddComponent<MeshFilter>();
            curtain.AddComponent<MeshRenderer>().sharedMaterial = sphere.GetComponent<MeshRenderer>().sharedMaterial;
            _curtain = curtain.AddComponent<DrapeCloth>();
            _curtain.Columns = 48;
            _curtain.Rows = 48;
            _curtain.Size = new Vector2(2f, 2f);
            _curtain.PinMode = DrapePinMode.None;
            _curtain.TotalMass = 0.4f;
            _curtain.SleepThreshold = 0.01f;
            _curtain.SleepTime = 1f;
            _curtain.PauseWhenInvisible = false;
            _curtain.Colliders.Colliders.Add(sphere.GetComponent<SphereCollider>());
            _curtain.Colliders.Planes.Add(floor.transform);
            _curtain.Colliders.Margin = 0.01f;
            _curtain.Colliders.Friction = 0.6f;
            curtain.SetActive(true);
            _nextDrop = Time.time + DropEvery;

            SampleSetup.CameraAndLight(new Vector3(0f, 2.5f, -4f), new Vector3(0f, 0.8f, 0f));
        }

        private void Update()
        {
            if (_curtain == null || DropEvery <= 0f || Time.time < _nextDrop) return;
            _nextDrop = Time.time + DropEvery;
            // Disabling releases the native cloth; enabling builds it again at its start pose.
            _curtain.enabled = false;
            _curtain.enabled = true;
        }
    }
}
